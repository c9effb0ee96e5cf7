"""jackpy.body"""
