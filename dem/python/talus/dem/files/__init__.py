"""Files in and out: checkpoints (and which may run Python), ParaView output, text export and import, mesh import."""
