"""tricycle"""
