"""The checks along a program: reach, joint limits and motors (motion.py), the gun body's
clearance from the part (clearance.py) and a cell's robots' from each other and the part
(cell_clearance.py), and what the drives' compliance does to the paint (compliance.py,
cell_compliance.py) (docs/model.md §21, §25, §26.4, §27.7)."""

# Nothing imported here: the planners below the kinds import single checks (line.panel the
# clearance), and compliance.py reads the planners' plans, so importing it here is a cycle.
# Each check is public in its module (compliance.program_deflection, compliance_entry, …).
__all__: list[str] = []
