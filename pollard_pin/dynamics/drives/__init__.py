"""The drives as springs (docs/model.md §27, §28): the static stiffness, deflection and modes
of compliant drives on rigid links, and the flexible-joint simulation's drives and plant."""
