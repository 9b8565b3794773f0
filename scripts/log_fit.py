"""The least-squares line a + b·log10 N through the permanent settlement after N load
cycles: what fig_cycles.py draws through the replicates' mean and what compare.py
reports per decade of cycles (b, the settlement per decade)."""
import numpy as np


def log_fit(cycles, settlement):
    """(a, b) of the least-squares line settlement = a + b·log10 N."""
    b, a = np.polyfit(np.log10(np.asarray(cycles, dtype=float)), settlement, 1)
    return a, b
