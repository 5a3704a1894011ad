"""AIS input: NMEA and CSV decoding, track cleaning, tracks written to bags."""
