"""Seed genetic algorithm over float gene arrays (ask/tell), its operators, seeds and seed pool."""
