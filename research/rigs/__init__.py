"""Study rigs: simulated experiments that the research scripts and the tests run, not the
levels the package ships.

- :mod:`research.rigs.pickup`: a roller picking chain up from a table or putting it down
  (the paper's section "Pick-Up and Pull-Down Forces"), alone in its own pymunk space.
- :mod:`research.rigs.cart_step`: a step in the upper cart's force on ``apparatus_floor``,
  measured against the energy balance (:func:`chainfountain.theory.apparatus.cart_step_speed`).
"""
