// Module tfm: filled in by its issue.
