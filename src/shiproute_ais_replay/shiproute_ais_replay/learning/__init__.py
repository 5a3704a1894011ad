"""Learning a ship model from its own records: records in (bags, CSV logs) with met along the
track, ISO 19030-style cleaning, synthetic records of a fouled ship, drift, CLI and bench."""
