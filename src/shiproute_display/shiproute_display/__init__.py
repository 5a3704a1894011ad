"""The bridge display: a live web page of plan, ship and forecast, and Foxglove topics."""
