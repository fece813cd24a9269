"""The analytic layer, numpy only (docs/model.md §7): ``closed_form`` (the thesis' IK with exact
jet derivatives), ``jet`` (forward-mode Taylor jets), ``taskspace`` (pose conventions).
Kept import-free so that it never pulls in Pinocchio."""
