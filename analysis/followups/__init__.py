"""Room 6, the follow-ups of an omnibus effect.

``paired`` (a paired difference), ``simple_effects`` (each factor within the levels of the others), ``pairwise``
(paired comparisons of levels), and for mixed designs ``pooled_followups`` (the pooled within-group covariance, as
emmeans on afex) and ``mixed_followups`` (which also keeps the per-group error). Imports only earlier rooms.
"""
