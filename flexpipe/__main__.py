from flexpipe.cli import main

raise SystemExit(main())
