"""Studies across models: the small-angle models against "paper" (:mod:`.compare`), every
model against the engines (:mod:`.validation`), and the built-in example (:mod:`.demo`)."""
