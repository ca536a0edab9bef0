"""The columns of the long table every input becomes (one definition for the package)."""

#: The long table's columns: ids (text), time t (s), positions x, y, z (m, the book's frame) and contact.
COLUMNS = ("participant", "trial", "t", "x", "y", "z", "contact")
ID_COLUMNS = ("participant", "trial")  #: the columns naming a trial (text)
POSITION_COLUMNS = ("x", "y", "z")  #: the position columns (m; y vertical)
