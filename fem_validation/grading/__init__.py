"""Graders: a result (ours or another code's) against Hertz.  They
never import a source."""
