Diagram s
  type Symmetrical
  theta 3
  phi 2
  NormalFlux 5
  def
  1 2 3
  4 5 6
enddef
Light a
  type area
  TotalFlux 5
  Diagram s
enddef
Fixture x
  Light a
  Position 0 0 0
  Direction 0 0 0
enddef
Group g
  Switch off
  def
  x
enddef
