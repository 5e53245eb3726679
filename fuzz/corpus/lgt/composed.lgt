Diagram c
  type AxiSymmetrical
  theta 4
  phi 1
  diagrams 2

  angle 30.00
  NormalFlux 100.0
  def
    10 5 1 0
  angle 60.00
  NormalFlux 100.0
  def
    8 6 2 0
enddef
Light L
  TotalFlux 10
  SpotLight on
  Diagram c
enddef
Fixture F
  Light L
  Position 0 1 0
enddef
