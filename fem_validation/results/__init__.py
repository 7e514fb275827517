"""What every source produces and every grader reads: one contact result
type (:mod:`.contact`) and one tangential one (:mod:`.tangential`)."""
