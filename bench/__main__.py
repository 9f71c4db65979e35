"""`python -m bench SUBCOMMAND ...` from a checkout: the same as `termpool bench SUBCOMMAND ...`."""

from bench import main

raise SystemExit(main())
