"""Cube-4 reports, apart from the simulation: ``gates`` (Yosys gate count per unit),
``fpga`` (ECP5 synthesis, place and route), ``report`` (image error against run time);
``synth`` is the synthesis plumbing the first two share, ``markdown`` the tables and the
provenance stamp (git commit, RTL digest) all of them write. Run them as
``python -m cube4_reports.<name>`` (``make gates``, ``make fpga``, ``make report``).
"""
