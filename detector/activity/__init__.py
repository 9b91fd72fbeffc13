"""Seed 001's nine (in)activity detectors (Olivares et al., "Detection of (In)activity Periods in Human
Body Motion Using Inertial Sensors: A Comparative Study", section 2), batch and streaming.

``common`` (the shared interface: ActivityResult, input checks, the sliding-window stream),
``magnitude`` (AMVD, AMD, ARED, SHOD, FRD: section 2.1), ``spectrum`` (LTSD, FSD: section 2.2),
``memory`` (MBGTD, MBCD: section 2.3) and ``registry`` (name -> detector). Nothing is imported here.
"""
