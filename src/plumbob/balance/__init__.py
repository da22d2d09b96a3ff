"""Make it stand: what to change so a body meets a stability target.

(This branch's placeholder: the balance room's own ``__init__`` exports its
public names; hollowing is :mod:`plumbob.balance.hollow`.)
"""
