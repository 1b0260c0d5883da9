"""Files: reading user files within bounds, atomic writes, output targets.

``files.py`` reads a user's file safely (regular files only, never past a limit), writes
and fsyncs bytes, and locks folders; ``journal.py`` is the record that makes a set of
files all-or-nothing across a kill; ``targets.py`` checks an output path before anything
is rendered, tells a file scanplan wrote from one it did not, and locks the output
folders; ``atomic.py`` writes one file or a set of files as a transaction. Each imports
only those before it. ``kept.py`` is the bounded memory every layer keeps what a re-plan
asks again in.
"""
