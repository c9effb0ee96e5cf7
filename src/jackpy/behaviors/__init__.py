"""jackpy.behaviors"""
