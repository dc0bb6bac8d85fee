import sys

from dynstiff.cli import main

sys.exit(main())
