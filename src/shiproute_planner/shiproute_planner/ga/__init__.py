"""Generic genetic algorithm over float gene arrays (ask/tell): operators, ranking, islands and
the seed pool. Knows nothing of routes: problems come in as bounds, arrays and callables."""
