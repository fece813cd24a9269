"""Shipped model description: parameters (TOML), URDF and SRDF (installed as pollard_pin.models)."""
