"""One run: the pipeline (fly -> sense -> detect -> path -> write, :mod:`.pipeline`), the run folder's
files (:mod:`.run_io`) and the recording's view of a run (:mod:`.run_view`)."""
