"""jackpy.analysis"""
