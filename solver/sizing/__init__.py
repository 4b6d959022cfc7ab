"""Sizing loads: the certification rules' load factors and design speeds (regulations), the gust
load factors of CS-23.341 (gusts), and the V-n diagram with the load cases it gives (vn, cases)."""
