"""The science, pure and fast: world rules, layouts, FOV, knowledge base, human model, belief, planners.

No I/O, no web, no database: everything here is a function of its arguments (randomness included,
through a ``numpy.random.Generator`` passed in).
"""
