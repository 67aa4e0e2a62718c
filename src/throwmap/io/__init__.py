"""Files: part/arm config files in TOML or JSON (:mod:`.config`), atomic writes and strict
JSON (:mod:`.files`)."""
