"""``yade._customConverters``: in Yade, the C++ module that registers Python <-> C++ converters
for its containers. Talus's bindings convert on their own, so the module is empty and
``from yade._customConverters import *`` (Yade's test modules start with it) imports nothing."""

__all__: list[str] = []
