"""What the solver can be asked: one input type per operation, each holding everything its
answer depends on and answering itself with `run()` (what a worker runs), and the one table of
operations (`table`) the web service derives its routes, jobs and documentation from.
"""
