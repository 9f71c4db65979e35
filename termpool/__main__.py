from termpool.cli import main

raise SystemExit(main())
