// Module coupling: filled in by its issue.
