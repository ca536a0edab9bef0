"""The paper's clustering settings, in a module that imports nothing (the command line reads them)."""

DEFAULT_K = 6  #: the paper's number of clusters (Sect. 6)
