"""The package's version: a leaf, so that any layer can stamp its outputs without importing the
package root."""
__version__ = "0.1.0"
