"""The model layer: parameters (TOML), the URDF/SRDF generator and the Pinocchio model with its
two cut spherical joints (docs/model.md §3–§5). Import the modules: ``params``, ``urdf``,
``build``. (Kept import-free so that numpy-only users never load Pinocchio.)"""
