// Module io: filled in by its issue.
