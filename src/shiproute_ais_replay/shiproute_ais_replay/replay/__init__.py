"""Voyage replay: bag messages scheduled on the bag clock at a chosen rate."""
