"""The command line: argument parsing and exit statuses only, one module
a mode (:mod:`.common` holds what they share)."""
