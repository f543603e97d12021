"""``python -m ironbark_opt.cli``: the ``ironbark`` command."""
from ironbark_opt.cli import main

main()
