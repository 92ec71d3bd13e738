"""Measurements and reports of a run: Yade's measures, energy, timing, progress, reference solutions and sliding-block experiments."""
