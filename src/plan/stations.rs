//! Truck stations: splitting a message so every stroke is reachable from one station.
