"""Fleet triage (`hexar triage`): every task of every recording under some folders, explained without an LLM.

inputs: which recordings the arguments name, and a label for each; work: one recording's rows, the unit of work
the runners hand out; local: a process pool; on_ray: Ray; command: the resumable run and its results file;
report: the tables, Markdown report and figures; compare: two runs or periods side by side.
"""
