"""Bad-input corpus: generators ``gen_*.py`` and the runner that loads every case."""
