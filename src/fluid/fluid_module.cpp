// Module fluid: filled in by its issue.
