"""Physically impossible forecast values: the limits ingest masks and validation refuses.

Limits (beyond any sea or atmosphere on record, so only decoding faults and fill values that
were not declared reach them): significant wave heights above 30 m or below 0 (the largest
measured Hs is ~19 m, WMO 2016; the largest modelled in hurricanes ~ 20 m), 10 m wind speeds
above 100 m/s (the strongest measured gust is 113 m/s, sustained winds stay below ~ 90 m/s),
wave periods <= 0 s or above 40 s (ocean wind waves and swell: 1-30 s), surface current speeds
above 5 m/s (the Gulf Stream, Kuroshio and Agulhas peak at 2.5-3 m/s), and infinities
anywhere.
"""

from __future__ import annotations

HS_MAX_M = 30.0
WIND_SPEED_MAX_M_S = 100.0
PERIOD_MAX_S = 40.0
CURRENT_SPEED_MAX_M_S = 5.0
