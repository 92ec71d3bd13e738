"""Controllers: time steppers, stress/strain controllers, triaxial engines, Peri3d, PID servo, Yade's scene generators."""
