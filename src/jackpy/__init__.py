"""jackpy: an interactive workbench for articulated human figures, after Penn's Jack."""

__version__ = "0.1.0"
