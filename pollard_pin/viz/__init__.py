"""What people look at: ``viewer`` (MeshCat, static HTML), ``plots`` (matplotlib figures) and
``report`` (sizing table and cross-checks)."""
