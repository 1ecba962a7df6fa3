# Independent bound on the first frequency of example 09 (README "Natural frequencies"):
# the links made rigid, a Rayleigh-Ritz subspace of the beam model (numpy).
import numpy as np
pi=np.pi
def tube(d,t): di=d-2*t; return pi*(d**2-di**2)/4, pi*(d**4-di**4)/64
Al,St=2700,7850
A1,I1=tube(0.1,0.005); A2,I2=tube(0.08,0.004); A3,I3=pi*0.04**2/4, pi*0.04**4/64
links=[(0,0.6,Al,A1,I1,1),(0.6,1.1,Al,A2,I2,2),(1.1,1.25,St,A3,I3,3)]
piv=[0.0,0.0,0.6,1.1]
def vel(x,b):
    c=np.zeros(4)
    for k in range(b+1): c[k]=x-piv[k]
    return c
def rot(b):
    c=np.zeros(4); c[:b+1]=1; return c
M=np.zeros((4,4))
xs,ws=np.polynomial.legendre.leggauss(6)
for x0,x1,rho,A,I,b in links:
    for xi,wi in zip(xs,ws):
        x=x0+(x1-x0)*(xi+1)/2; w=wi*(x1-x0)/2
        c=vel(x,b); M+=rho*A*w*np.outer(c,c)
    r=rot(b); M+=rho*I*(x1-x0)*np.outer(r,r)
for m,Iyy,x,b in [(6,0.03,0.6,1),(3,0.008,1.1,2)]:
    c=vel(x,b); M+=m*np.outer(c,c); r=rot(b); M+=Iyy*np.outer(r,r)
Ac,Ic=tube(0.14,0.008); L=0.5
mc=0
for xi,wi in zip(xs,ws):
    s=(xi+1)/2; w=wi*L/2
    mc+=Al*Ac*w*(L*(s**3-s**2))**2 + Al*Ic*w*(3*s**2-2*s)**2
M[0,0]+=mc
E=70e9; kc=4*E*Ic/L
K=np.diag([kc,2e5,1e5,3e4])
ev=np.sort(np.linalg.eigvals(np.linalg.solve(M,K)).real)
print("kc %.4g  f (Hz):"%kc,np.sqrt(ev)/2/pi)
ev2=np.sort(np.linalg.eigvals(np.linalg.solve(M[1:,1:],K[1:,1:])).real); print("rigid column:",np.sqrt(ev2)/2/pi)
