"""Studies over many flights: the detector sweep (:mod:`.sweep`), certification (:mod:`.certify`) and
the checks of a run or a population against public anchors (:mod:`.validate`)."""
