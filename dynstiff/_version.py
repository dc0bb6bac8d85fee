"""The package's version (read by the command line, the reports and the metadata of every
file written)."""

__version__ = "0.1.0"
