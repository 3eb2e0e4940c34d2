"""The command line's commands, one module per capability; :mod:`amiro.cli` builds the parser.

Each module keeps its heavy imports inside its handlers, so `amiro --help` answers at once."""
