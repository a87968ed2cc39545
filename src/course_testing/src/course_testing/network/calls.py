#!/usr/bin/env python3
"""Make service calls from one process and print, as one JSON list, what each call returned.

    calls.py '[["/spawn", {"name": "a b", "x": 1.0}], ...]'

Each result is {"ok": true, "response": {field: value}} or {"ok": false, "error": text}; fields the
service does not have fail on the client side with the error a user would read from rosservice.
"""
import json
import sys

import rospy
import rosservice


def call(service, fields):
    try:
        service_class = rosservice.get_service_class_by_name(service)
        response = rospy.ServiceProxy(service, service_class)(**fields)
    except (rospy.ServiceException, rosservice.ROSServiceException, TypeError, ValueError) as error:
        return {'ok': False, 'error': str(error)}
    return {'ok': True, 'response': {slot: getattr(response, slot) for slot in response.__slots__}}


def main():
    rospy.init_node('calls', anonymous=True, disable_signals=True)
    results = [call(service, fields) for service, fields in json.loads(sys.argv[1])]
    print(json.dumps(results), flush=True)


if __name__ == '__main__':
    main()
