/**
 * Bus members that the tests start in JVMs of their own. They live outside
 * {@code io.dtron.api} so that they can use nothing but its public API.
 */
package io.dtron.testadapter;
