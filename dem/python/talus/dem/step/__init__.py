"""The engines of a time step with Yade's names: the core engines, Python engines, force and kinematic engines, the domain limiter, Yade's older spellings."""
