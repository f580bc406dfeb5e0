"""``python -m viscosine`` and the ``viscosine`` command: the command line of
``python -m comparisons`` (the same parser, `comparisons.cli`), under the name it was called by."""
import sys

from comparisons import cli


def main(argv=None):
    """The ``viscosine`` console script: run the command line, return its exit status."""
    return cli.main(argv, prog="viscosine")


if __name__ == "__main__":
    sys.exit(cli.main(prog="python -m viscosine"))
