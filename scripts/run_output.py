"""Reading an estep run's history.csv for the figure scripts, with one clear message.

read_history() ends the script (exit status 1) with a line naming the file and what is wrong
with it, before the script draws anything: a file it cannot read, one without rows, one without
a column the figure needs (the history of another problem), or a row that is not numbers (a
file cut short).
"""
import csv
import os
import sys


def fail(message):
    """End the calling script with `<script>: error: message` and exit status 1."""
    sys.exit(f"{os.path.basename(sys.argv[0])}: error: {message}")


def read_history(path, columns):
    """The history file at path as {column: list of floats}; it must hold the given columns."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as error:
        fail(f"cannot read <{path}>: {error.strerror}")
    if not rows:
        fail(f"<{path}> has no rows")
    missing = [c for c in columns if c not in rows[0]]
    if missing:
        fail(f"<{path}> has no column {', '.join(missing)}: is it the history of the run "
             "this figure draws?")
    # The header ends with a comma: its last, empty name is no column.
    history = {key: [] for key in rows[0] if key}
    for line, row in enumerate(rows, start=2):
        for key, values in history.items():
            try:
                values.append(float(row[key]))
            except (TypeError, ValueError):
                fail(f"<{path}>, line {line}: column {key} holds <{row[key]}>, not a number "
                     "(a file cut short?)")
    return history
