;; written for raygine's fuzz corpus

Geography Somewhere
  zenith    0.0000 1.0000 0.0000
  latitude  48.0
  time      09:30
enddef

Diagram down
  type AxiSymmetrical
  theta  7
  phi   1
  NormalFlux 1000.0000
  def
    300.0 280.0 220.0 120.0 40.0
    0.0 0.0
enddef

Light Lp
  type point
  TotalFlux  1200.0000
  intensity  1.0000 0.9000 0.8000
  heat off
  CastShadows on
  SpotLight  off
enddef

Light Ld
  type point
  TotalFlux  800.0
  intensity  1 1 1
  Diagram down
enddef

Fixture F1
  Light   Lp
  Switch  on
  GeLight off
  Position  1.0 2.5 -1.0
  Direction 0.0000 -1.0000 0.0000
  Rotation  0.0000
enddef

Fixture F2
  Light   Ld
  Switch  on
  Position  3.0 2.5 -1.0
  Direction 0.0 -1.0 0.0
  Rotation  30.0
enddef

Fixture F3
  Light   Lp
  Switch  off
  Position  2.0 2.5 -3.0
enddef

Group main
  Switch on
  Edit   on
  Shown  on
  Power  75.0%
  def
    F1
    F2
    F3
enddef
