"""An example lab's robots for Steakhouse Study (README.md beside this package): ``mylab_scripted``, a robot that
follows a fixed recipe, and ``mylab_learned``, a policy over the same skills learned by Q-learning in the kitchen
environment (``train.py``)."""
