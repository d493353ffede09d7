"""Brushing policies (thesis chapter 3) that drive ``hairbrush_env``; this package may import
``hairbrush_env``, never the reverse."""
