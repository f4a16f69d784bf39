"""Screw-rotor profile families as rack chains (Rinder, *Sonderverzahnungen für Schraubenverdichterrotoren*, sec. 1.2)."""
