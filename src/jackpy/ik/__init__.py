"""jackpy.ik"""
