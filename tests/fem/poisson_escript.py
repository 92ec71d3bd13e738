"""The same Poisson problem with escript (finley, order 2), run by run-escript: the escript-style
driver of fem/ assembles LinearPDE objects like this one."""
from esys.escript import *
from esys.escript.linearPDEs import LinearPDE
from esys.finley import Rectangle
dom = Rectangle(8, 8, order=2)
x = dom.getX()
pde = LinearPDE(dom)
mask = whereZero(x[0]) + whereZero(x[0]-1) + whereZero(x[1]) + whereZero(x[1]-1)
exact = 1 + x[0]**2 + 2*x[1]**2
pde.setValue(A=kronecker(dom), Y=-6, q=mask, r=exact)
u = pde.getSolution()
print("err", Lsup(u - exact))
