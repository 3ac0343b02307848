"""``python -m spiralbevel``: the same command line as ``spiralbevel``."""

from .cli import main

if __name__ == "__main__":  # pragma: no branch
    main()
