"""jackpy.devices"""
