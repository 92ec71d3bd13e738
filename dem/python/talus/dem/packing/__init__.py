"""Packings and particle insertion: lattices and clouds clipped by predicates, dense random packings, factories, reset positions, moving groups of bodies."""
