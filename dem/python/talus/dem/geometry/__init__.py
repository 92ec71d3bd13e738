"""Shapes and boundary geometry: spheres, walls, facets, boxes, Potential Blocks and Particles, block generation, triangulated surfaces, how bodies look."""
