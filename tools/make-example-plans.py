# Writes the plans of examples/ (the gallery figures, docs/gallery.md). Geometry helpers below;
# each block names the mesh and the frame it is written in. python3 tools/make-example-plans.py
import json, math
import os
OUT=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'examples') + '/'
def sub(a,b): return [a[i]-b[i] for i in range(3)]
def add(a,b): return [a[i]+b[i] for i in range(3)]
def mul(a,s): return [x*s for x in a]
def dot(a,b): return sum(a[i]*b[i] for i in range(3))
def cross(a,b): return [a[1]*b[2]-a[2]*b[1],a[2]*b[0]-a[0]*b[2],a[0]*b[1]-a[1]*b[0]]
def nrm(a): n=math.sqrt(dot(a,a)); return mul(a,1/n)
def rot(v,k,ang):
    k=nrm(k); c,s=math.cos(ang),math.sin(ang)
    return add(add(mul(v,c),mul(cross(k,v),s)),mul(k,dot(k,v)*(1-c)))
def r(v,n=6): return [(round(x,n)+0.0 if abs(x-round(x,n))<1e-13 else x) for x in v]
def end(p,t,n): return {"position":r(p),"tangent":r(t),"normal":r(n)}
def ribbon(p0,t0,n0,p1,t1,n1,turns=0):
    d={"start":end(p0,t0,n0),"end":end(p1,t1,n1)}
    if turns: d["extraTurns"]=turns
    return d
def warp(ini,fin,R,shape="bell",p=None,sub=None,name=None):
    w={}
    if name: w["name"]=name
    w["initial"]=ini; w["final"]=fin; w["radius"]=R
    w["decay"]={"shape":shape} if shape=="bell" else {"shape":shape,"plateau":p}
    if sub: w["subdivision"]={"tolerance":sub[0],"maxPasses":sub[1]}
    return w
def plan(fn,name,warps,units="mm"):
    d={"format":"bender-warps","version":1,"units":units,"name":name,"warps":warps}
    s=json.dumps(d,indent=2)
    # keep the short vectors on one line
    import re
    s=re.sub(r'\[\s+([-0-9.e]+),\s+([-0-9.e]+),\s+([-0-9.e]+)\s+\]',r'[\1, \2, \3]',s)
    open(OUT+fn,'w').write(s+'\n')
def bend(p0,t,n_bend_axis,L,phi,u):
    """Arc of length L starting at p0 with tangent t turning by phi towards u."""
    if phi==0: return add(p0,mul(t,L)),t
    rho=L/phi
    return add(p0,add(mul(t,rho*math.sin(phi)),mul(u,rho*(1-math.cos(phi))))), add(mul(t,math.cos(phi)),mul(u,math.sin(phi)))
def straight(p0,t,n,L): return ribbon(p0,t,n,add(p0,mul(t,L)),t,n)

# --- display helper: y-up meshes (CGAL data) to z-up for bender-cli render, a rigid warp
X=[1,0,0]
plan('display-y-up-to-z-up.bender.json',
  'display helper: rotate a y-up mesh by 90 degrees about x (y -> z); rigid: the plateau covers everything',
  [warp(straight([-1,0,0],X,[0,0,1],2), straight([-1,0,0],X,[0,-1,0],2), 100.0,'plateau',0.95)],units='model')

# --- Fig. 1: the cow (y up, head +x, legs -y, lateral z)
Y=[0,1,0]; mY=[0,-1,0]; Z=[0,0,1]
W=[]
def legs(x, fwd, name, phi):
    p0=[x,-0.09,0]; L=0.24
    p1,t1=bend(p0,mY,Z,L,phi,[fwd,0,0])
    return warp(ribbon(p0,mY,Z,add(p0,mul(mY,L)),mY,Z), ribbon(p0,mY,Z,p1,t1,Z),0.17,'plateau',0.75,name=name)
W.append(legs(0.13, 1, 'front legs bent forwards', math.radians(75)))
W.append(legs(-0.355,-1, 'hind legs bent backwards', math.radians(70)))
for sz in (1,-1):
    b=[0.33,0.283,0.045*sz]; tip=[0.42,0.31,0.08*sz]; L=math.dist(b,tip)*1.15
    t=nrm(sub(tip,b)); n=nrm(cross(t,[0,0,1]))  # normal in the horn's vertical plane
    dv=[0,-1,0.9*sz]
    down=nrm(sub(dv,mul(t,dot(dv,t))))
    p1,t1=bend(b,t,None,L,math.radians(75),down)
    n1=nrm(cross(t1,cross(n,t)))  # keep the bending axis
    n0=nrm(cross(cross(t,n),t)) if False else n
    ax=nrm(cross(t,down)); n0=nrm(cross(ax,t)); n1=nrm(cross(ax,t1))
    W.append(warp(ribbon(b,t,n0,add(b,mul(t,L)),t,n0), ribbon(b,t,n0,p1,t1,n1),0.035,'plateau',0.6,
      name='%s horn bent downwards'%('left' if sz>0 else 'right')))
# humps: the back, an S-shaped wire with the same ends
p0=[-0.38,0.16,0]; p1=[0.08,0.16,0]; tt=nrm([1,1.1,0])
W.append(warp(ribbon(p0,X,Y,p1,X,Y), ribbon(p0,tt,nrm(cross(Z,tt)),p1,tt,nrm(cross(Z,tt))),0.15,'bell',name='humps on the back'))
# neck: stretched forwards; the head moves rigidly inside the plateau
p0=[0.12,0.1,0]; t=nrm([1,0.6,0]); n=nrm(cross(Z,t)); L=0.2
W.append(warp(ribbon(p0,t,n,add(p0,mul(t,L)),t,n), ribbon(p0,t,n,add(p0,mul(t,L+0.08)),t,n),0.3,'plateau',0.75,name='neck stretched'))
plan('fig01-cow.bender.json','Fig. 1: the cow in 6 warps (legs, horns, humps, neck)',W,units='model')

# --- Fig. 2: the bunny's ear (bunny00.off: y up; the upright ear, wide along x)
b=[-0.08,0.335,-0.03]; tip=[-0.01,0.5,-0.118]; L=math.dist(b,tip)
t=nrm(sub(tip,b)); wdir=[1,0,0]; n=nrm(cross(t,wdir))
ax=wdir  # bend about the ear's width direction
u=nrm(cross(ax,t))
p1,t1=bend(b,t,None,L,math.radians(60),u)
n1=nrm(cross(t1,ax))
ini=ribbon(b,t,n,add(b,mul(t,L)),t,n)
bentR=ribbon(b,t,n,p1,t1,n1)
bendW=warp(ini,bentR,0.13,'plateau',0.5,name='ear bent')
plan('fig02-bunny-ear-bend.bender.json','Fig. 2: the bunny ear bent',[bendW],units='model')
# then twisted: grab the bent ear again and turn its tip by 120 degrees about the wire
n1t=rot(n1,t1,math.radians(90))
twistW=warp(bentR, ribbon(b,t,n,p1,t1,n1t),0.1,'plateau',0.5,name='ear twisted')
plan('fig02-bunny-ear-bend-twist.bender.json','Fig. 2: the bunny ear bent, then twisted',[bendW,twistW],units='model')

# --- Fig. 8: unit-diameter sphere (sphere.off, radius 0.5) grabbed by a nearly closed circle
rho=0.5; g=0.025
ini={"start":end([rho*math.cos(g),rho*math.sin(g),0],[-math.sin(g),math.cos(g),0],Z),
     "end":end([rho*math.cos(g),-rho*math.sin(g),0],[math.sin(g),math.cos(g),0],Z)}
fin=ribbon([-0.25,0.75,0],[-1,0,0],Z,[-0.25,-0.75,0],[1,0,0],Z)
plan('fig08-sphere-circle.bender.json','Fig. 8: a sphere grabbed by a nearly closed circle that opens',
  [warp(ini,fin,0.25,'bell')],units='model')

# --- Tube (tests/data/conformance/tube.off): axis x from 0 to 40, radius 5, y, z lateral
ZZ=[0,0,1]; YY=[0,1,0]
def tubeplan(fn,name,fin,p0=[20,0,0],L=20,R=8,shape='plateau',p=0.75,sub=None,ini=None):
    ini=ini or straight(p0,X,YY,L)
    plan(fn,name,[warp(ini,fin,R,shape,p,sub)])
# Fig. 9: a rigid motion of the wire: bell vs plateau (the tube spans x in [-5, 45])
O9=[25,0,0]
G=lambda v: add(rot(sub(v,O9),YY,math.radians(-50)),[0,0,6])
G=(lambda g: (lambda v: add(g(v),O9)))(G)
Gv=lambda v: rot(v,YY,math.radians(-50))
fin9=ribbon(G([25,0,0]),Gv(X),Gv(YY),G([47,0,0]),Gv(X),Gv(YY))
tubeplan('fig09-tube-bell.bender.json','Fig. 9: rigid motion of the wire, bell decay',fin9,p0=O9,L=22,shape='bell')
tubeplan('fig09-tube-plateau.bender.json','Fig. 9: rigid motion of the wire, plateau decay',fin9,p0=O9,L=22,shape='plateau',p=0.75)
# Fig. 10: the tip turned 200 degrees about the wire: the minimal screw flips at s = 0.9
p1,t1=bend([5,0,0],X,None,42,math.radians(90),ZZ)
tubeplan('fig10-tube-flip.bender.json','Fig. 10: bend of 90 degrees with a twist of 200 degrees (the minimal screw axis flips)',
  ribbon([5,0,0],X,YY,p1,t1,rot(YY,t1,math.radians(200)),turns=1),p0=[5,0,0],L=42,R=8,shape='bell')
# Fig. 14 (wires run past the tube's end at x = 45 so that the end moves with them)
p1,t1=bend([25,0,0],X,None,22,math.radians(90),ZZ)
tubeplan('fig14-tube-bend.bender.json','Fig. 14: bend',ribbon([25,0,0],X,YY,p1,t1,YY),p0=[25,0,0],L=22)
tubeplan('fig14-tube-twist.bender.json','Fig. 14: twist',
  ribbon([-7,0,0],X,rot(YY,X,math.radians(-150)),[47,0,0],X,rot(YY,X,math.radians(150))),p0=[-7,0,0],L=54)
tubeplan('fig14-tube-stretch.bender.json','Fig. 14: stretch',ribbon([10,0,0],X,YY,[60,0,0],X,YY),p0=[10,0,0],L=37)
th=math.radians(250)
p1,t1=bend([5,0,0],X,None,42,th,ZZ)
tubeplan('fig14-tube-curl.bender.json','Fig. 14: curl',ribbon([5,0,0],X,YY,p1,t1,YY),p0=[5,0,0],L=42,R=6.5,p=0.8)
p1,t1=bend([27,0,0],X,None,20*1.3,math.radians(180),ZZ)
tubeplan('fig14-tube-hook.bender.json','Fig. 14: hook',ribbon([27,0,0],X,YY,p1,t1,YY),p0=[27,0,0],L=20,R=6.5,p=0.8)

# --- Fig. 13 and 11: plane.off (y = 0, x and z in [-0.625, 0.625]); subdivision refines
SUB=(0.002,6)
def pplan(fn,name,ini,fin,R,shape='bell',p=None,sub=SUB):
    plan(fn,name,[warp(ini,fin,R,shape,p,sub)],units='model')
# bowl: a short wire through the plane, pushed down
pplan('fig13-plane-bowl.bender.json','Fig. 13: bowl',straight([0,-0.1,0],Y,X,0.2),straight([0,-0.4,0],Y,X,0.2),0.55,'plateau',0.25)
# wave: a straight wire along x turned into an S
tt=nrm([1,1.2,0])
pplan('fig13-plane-wave.bender.json','Fig. 13: wave',straight([-0.6,0,0],X,Y,1.2),
  ribbon([-0.6,0,0],tt,nrm(cross(ZZ,tt)),[0.6,0,0],tt,nrm(cross(ZZ,tt))),0.5)
# fin: a straight wire along x lifted
pplan('fig13-plane-fin.bender.json','Fig. 13: fin',straight([-0.35,0,0],X,Y,0.7),straight([-0.35,0.3,0],X,Y,0.7),0.16)
# embossed S: an S-shaped wire (two semicircles) raised
Sini=ribbon([0,0,-0.36],X,Y,[0,0,0.36],X,Y)
Sfin=ribbon([0,0.05,-0.36],X,Y,[0,0.05,0.36],X,Y)
pplan('fig13-plane-emboss-s.bender.json','Fig. 13: embossed S',Sini,Sfin,0.07)
# horn: a wire ending just under the plane; its free end is pulled up and curled
p0=[0,-0.25,0]; ini=straight(p0,Y,X,0.24)
hp1,ht1=bend([0,-0.01,0],Y,None,0.6,math.radians(100),X)
pplan('fig13-plane-horn.bender.json','Fig. 13: horn',ini,ribbon(p0,Y,X,hp1,ht1,nrm(cross(ht1,ZZ))),0.3)
pplan('fig11-plane-horn-coarse.bender.json','Fig. 11: the horn on the original triangulation',ini,
  ribbon(p0,Y,X,hp1,ht1,nrm(cross(ht1,ZZ))),0.3,sub=None)

# --- Fig. 12: the aneurysm's widest vessel (aneurysm_data.stl, mm), its open end bent
P0=[12.4,-6.8,30.5]; Pend=[10.1,-24.6,39.4]; t=nrm(sub(Pend,P0)); L=math.dist(P0,Pend)+1.5
away=[2.8,3.5,7.6]; u=nrm(sub(away,mul(t,dot(away,t)))); ax=nrm(cross(t,u))
p1,t1=bend(P0,t,None,L,math.radians(60),u)
plan('fig12-aneurysm-bend.bender.json','Fig. 12: the aneurysm junction, one vessel bent',
  [warp(ribbon(P0,t,ax,add(P0,mul(t,L)),t,ax),ribbon(P0,t,ax,p1,t1,ax),7.0,'plateau',0.75)])
