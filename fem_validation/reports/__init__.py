"""Report writers: tables, figures and grade files from results and
grades handed to them (they import no solver and no run)."""
