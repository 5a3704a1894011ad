"""Route encoding (heading + RPM genes), generation stage by stage, evaluation and constraints."""
