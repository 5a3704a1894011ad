"""Geography: GSHHG land mask, geodesy helpers in a continuous longitude frame, port gazetteer."""
